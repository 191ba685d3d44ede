// Entry point: the debug object, the view registry and the router.
//
// To add a view, register its path with a function that mounts it and returns { unmount() }:
//   router.register( '/workbench', async ( container ) => ( await import( './ui/Workbench.js' ) ).mount( container ) );
// and link to it as `#/workbench`.

import './styles.css';
import './ui/nav.css';
import { installDebug, registerDebug } from './debug.js';
import { Router } from './ui/router.js';
import { NavBar } from './ui/NavBar.js';

installDebug( window );

// The navigation between the views: its own row above the views' container, never inside it.
const nav = new NavBar( { win: window } );
document.body.classList.add( 'has-nav' );
document.body.prepend( nav.element );
nav.start();

const router = new Router( document.getElementById( 'app' ) );

router.register( '/', async ( container ) => ( await import( './ui/HeadView.js' ) ).mountHeadView( container ), { title: 'Glasshead' } );
router.register( '/workbench', async ( container ) => ( await import( './ui/WorkbenchView.js' ) ).mountWorkbenchView( container ), { title: 'Glasshead workbench' } );
router.register( '/clinician', async ( container ) => ( await import( './ui/ClinicianView.js' ) ).mountClinicianView( container ), { title: 'Glasshead clinician' } );
router.register( '/speak', async ( container ) => ( await import( './ui/SpeechView.js' ) ).mountSpeechView( container ), { title: 'Glasshead: say it' } );
router.register( '/signin', async ( container ) => ( await import( './ui/SignInView.js' ) ).mountSignInView( container ), { title: 'Glasshead: sign in' } );
router.register( '/teach', async ( container ) => ( await import( './ui/LessonRunner.js' ) ).mountLessonRunner( container ), { title: 'Glasshead: lessons' } );
router.register( '/practice', async ( container ) => ( await import( './ui/ChildPractice.js' ) ).mountChildPractice( container ), { title: 'Glasshead: practise' } );
router.register( '/author', async ( container ) => ( await import( './ui/LessonEditor.js' ) ).mountLessonEditor( container ), { title: 'Glasshead: write lessons' } );
router.register( '/admin', async ( container ) => ( await import( './ui/AdminView.js' ) ).mountAdminView( container ), { title: 'Glasshead: privacy' } );

registerDebug( 'route', () => router.currentPath );
registerDebug( 'routes', () => router.paths );

router.start().catch( ( error ) => {

	console.error( 'Glasshead: the page could not start:', error );

} );

export { router };
