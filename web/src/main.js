// Entry point: the debug object, the view registry and the router.
//
// Each view has its folder under ui/ (head, workbench, speak, listen, clinician, lessons, practice,
// author, fits, admin, signin) with the modules only it uses; what two or more views use is in ui/shared. Every
// view extends ui/shared/View.js (mounting, clean-ups, the 3D stage) and loads through api.js.
// To add a view, register its path with a function that mounts it and returns { unmount() }:
//   router.register( '/workbench', async ( container ) => ( await import( './ui/workbench/WorkbenchView.js' ) ).mountWorkbenchView( container ) );
// and link to it as `#/workbench`.

import './styles.css';
import './ui/shared/nav.css';
import { installDebug, registerDebug } from './debug.js';
import { Router } from './ui/shared/router.js';
import { NavBar } from './ui/shared/NavBar.js';

installDebug( window );

// The navigation between the views: its own row above the views' container, never inside it.
const nav = new NavBar( { win: window } );
document.body.classList.add( 'has-nav' );
document.body.prepend( nav.element );
nav.start();

const router = new Router( document.getElementById( 'app' ) );

router.register( '/', async ( container ) => ( await import( './ui/head/HeadView.js' ) ).mountHeadView( container ), { title: 'Glasshead' } );
router.register( '/workbench', async ( container ) => ( await import( './ui/workbench/WorkbenchView.js' ) ).mountWorkbenchView( container ), { title: 'Glasshead workbench' } );
router.register( '/clinician', async ( container ) => ( await import( './ui/clinician/ClinicianView.js' ) ).mountClinicianView( container ), { title: 'Glasshead clinician' } );
router.register( '/speak', async ( container ) => ( await import( './ui/speak/SpeechView.js' ) ).mountSpeechView( container ), { title: 'Glasshead: say it' } );
router.register( '/signin', async ( container ) => ( await import( './ui/signin/SignInView.js' ) ).mountSignInView( container ), { title: 'Glasshead: sign in' } );
router.register( '/teach', async ( container ) => ( await import( './ui/lessons/LessonRunner.js' ) ).mountLessonRunner( container ), { title: 'Glasshead: lessons' } );
router.register( '/practice', async ( container ) => ( await import( './ui/practice/ChildPractice.js' ) ).mountChildPractice( container ), { title: 'Glasshead: practise' } );
router.register( '/author', async ( container ) => ( await import( './ui/author/LessonEditor.js' ) ).mountLessonEditor( container ), { title: 'Glasshead: write lessons' } );
router.register( '/listen', async ( container ) => ( await import( './ui/listen/ListenView.js' ) ).mountListenView( container ), { title: 'Glasshead: listen' } );
router.register( '/fits', async ( container ) => ( await import( './ui/fits/FitsView.js' ) ).mountFitsView( container ), { title: 'Glasshead: fit a target' } );
router.register( '/admin', async ( container ) => ( await import( './ui/admin/AdminView.js' ) ).mountAdminView( container ), { title: 'Glasshead: privacy' } );

registerDebug( 'route', () => router.currentPath );
registerDebug( 'routes', () => router.paths );

router.start().catch( ( error ) => {

	console.error( 'Glasshead: the page could not start:', error );

} );

export { router };
